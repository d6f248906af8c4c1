"""airfoil"""
