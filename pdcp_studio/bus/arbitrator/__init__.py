"""The bus arbitrator: pure deciders (claim, node table, presence) and its parts."""
