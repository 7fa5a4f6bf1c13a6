"""protocol tests"""
