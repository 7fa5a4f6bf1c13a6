"""The trace dock and its frame store, table models, captures and recording."""
