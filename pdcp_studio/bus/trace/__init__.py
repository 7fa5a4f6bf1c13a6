"""The trace: frame decoder, statistics, bus time, bulk transfers, what a listener learns;
capture files (formats, node map, replay) in ``files/``."""
