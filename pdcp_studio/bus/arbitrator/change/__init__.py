"""The change road on the bus: transactions and the interlock that holds devices still."""
