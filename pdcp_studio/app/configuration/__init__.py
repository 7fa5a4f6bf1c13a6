"""The window of one stored-configuration file (``.pdcfg``): its list, links and fit."""
