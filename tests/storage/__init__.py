"""storage tests"""
