"""The serial host link: the PC's client, the arbitrator's server, their records."""
