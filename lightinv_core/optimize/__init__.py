"""Optimisation: the design problem (F, G, penalty), the methods behind one run(problem,
context) and their registry.
"""
