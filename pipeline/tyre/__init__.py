"""tyre"""
