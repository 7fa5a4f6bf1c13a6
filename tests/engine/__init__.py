"""engine tests"""
