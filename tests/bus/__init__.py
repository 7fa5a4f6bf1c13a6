"""bus tests"""
