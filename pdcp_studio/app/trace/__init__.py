"""The trace dock and its frame store, table models, filters, search and markers; opening,
saving and recording captures in ``files/``."""
