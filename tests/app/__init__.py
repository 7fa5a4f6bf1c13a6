"""app tests"""
