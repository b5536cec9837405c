"""The inverse problem as data: sources, arrays, rules, intentions, goals, daylight;
variables, geometric rules, EN 12464-1 presets and solutions.
"""
