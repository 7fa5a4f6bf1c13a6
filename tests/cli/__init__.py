"""cli tests"""
