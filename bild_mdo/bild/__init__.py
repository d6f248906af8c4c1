"""bild"""
