"""Light transport by ray casting: form factors, reference radiosity solvers, photometric
luminaires, work planes, glazing under a sky.
"""
