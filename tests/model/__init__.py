"""model tests"""
