#!/usr/bin/python3
"""Write plate.csv, the particle file of the user guide's "check your own model":
a 0.2 m x 0.05 m plate, 41 x 11 particles 5 mm apart, the interior ones moved by up to
15% of the spacing in each direction (a user's particles are rarely a perfect lattice),
the left edge in group 'clamp', the others in group 'body'; no volume column (mfstab takes
the dual areas of the Delaunay triangulation).  usage: make_plate.py > plate.csv"""
import random

random.seed(15)
nx, ny, dx = 41, 11, 0.005
print("x,y,group")
for j in range(ny):
    for i in range(nx):
        x, y = i * dx, j * dx
        if 0 < i < nx - 1 and 0 < j < ny - 1:
            x += 0.15 * dx * (2 * random.random() - 1)
            y += 0.15 * dx * (2 * random.random() - 1)
        print(f"{x:.6f},{y:.6f},{'clamp' if i == 0 else 'body'}")
