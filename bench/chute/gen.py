#!/usr/bin/env python3
"""The granular chute of LAMMPS's benchmark inputs (bench/in.chute: 32,000
spheres of diameter 1 and density 1, a frozen rough base, Hooke law with
history k_n = 200000, gamma_n = 50 per unit m*, no tangential damping,
friction 0.5, gravity 1 tilted 26 degrees, dt = 1e-4, periodic in x and y)
as one set of initial positions for both codes: LAMMPS's data file is not
shipped with its Debian package, so the base and the bed are made here.

  gen.py WORK STEPS [NX] [LAYERS] [SEED] [ANGLE] [BASE]

writes WORK/data.chute and WORK/in.chute (LAMMPS) and WORK/case.yaml with
WORK/base.xyz and WORK/bed.xyz (grains). The base: NX x NX spheres on a
square lattice of spacing 1 in the plane z = 0, each moved by up to 0.3 in x
and y (a rough floor). The bed: LAYERS layers of NX x NX spheres on a
lattice of spacing 1.05 above it, each moved by up to 0.02 (no two touch).
ANGLE: the chute's inclination in degrees (default 26, LAMMPS's; the chute
flow case, cases/chute_flow, uses 24 as Silbert et al. 2001). BASE: lattice
(the default, as above) or random: NX x NX spheres at random positions no
closer than 0.7 in x and y, each at a random height in [-0.25, 0.25] (a
random rough floor, as Silbert et al.'s frozen random packing: a lattice
base lets a monodisperse flow order into layers), on a plane at z = 0 that
stops grains from falling through its gaps."""
import math
import random
import sys

work = sys.argv[1]
steps = int(sys.argv[2])
nx = int(sys.argv[3]) if len(sys.argv) > 3 else 40
layers = int(sys.argv[4]) if len(sys.argv) > 4 else 21
seed = int(sys.argv[5]) if len(sys.argv) > 5 else 1
angle = float(sys.argv[6]) if len(sys.argv) > 6 else 26.0
base_kind = sys.argv[7] if len(sys.argv) > 7 else "lattice"
end = "%.10g" % (steps * 1e-4)
rng = random.Random(seed)
L = float(nx)  # box side (base spacing 1)
if base_kind == "lattice":
    base = [((i + 0.5 + rng.uniform(-0.3, 0.3)) % L, (j + 0.5 + rng.uniform(-0.3, 0.3)) % L, 0.0)
            for i in range(nx) for j in range(nx)]
elif base_kind == "random":
    base = []
    while len(base) < nx * nx:  # random sequential addition, periodic in x and y
        x, y = rng.uniform(0, L), rng.uniform(0, L)
        if all(min(abs(x - p[0]), L - abs(x - p[0])) ** 2 + min(abs(y - p[1]), L - abs(y - p[1])) ** 2 >= 0.49
               for p in base):
            base.append((x, y, rng.uniform(-0.25, 0.25)))
else:
    sys.exit("gen.py: BASE is lattice or random, not " + base_kind)
z0 = 1.1 if base_kind == "lattice" else 1.35  # the bed's first layer clear of the base
s = L / math.floor(L / 1.05)  # bed spacing: a whole number of cells across the periodic box
m = int(round(L / s))
bed = []
for k in range(layers):
    for i in range(m):
        for j in range(m):
            bed.append(((i + 0.5) * s + rng.uniform(-0.02, 0.02), (j + 0.5) * s + rng.uniform(-0.02, 0.02),
                        z0 + k * s + rng.uniform(-0.02, 0.02)))
ztop = z0 + layers * s
zmax = ztop + 40.0

with open(work + "/base.xyz", "w") as f:
    for p in base:
        f.write("%.17g %.17g %.17g\n" % p)
with open(work + "/bed.xyz", "w") as f:
    for p in bed:
        f.write("%.17g %.17g %.17g\n" % p)

g = math.radians(angle)
floor = ("walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: grain}\n"
         if base_kind == "random" else "")
with open(work + "/case.yaml", "w") as f:
    f.write(f"""title: LAMMPS chute benchmark scene ({len(base) + len(bed)} spheres)
domain: {{min: [0, 0, -1], max: [{L}, {L}, {zmax}], periodic: [true, true, false]}}
gravity: [{math.sin(g):.17g}, 0, {-math.cos(g):.17g}]
materials:
  - {{name: grain, density: 1, youngs_modulus: 1e6, poisson_ratio: 0.3, restitution: 0.9, friction: 0.5}}
contact:
  model: linear
  tangential: linear
  linear: {{stiffness: 200000, damping_rate: 50, tangential_stiffness_ratio: 0.2857142857142857, tangential_damping_ratio: 0}}
particles:
  - {{name: base, material: grain, radius: 0.5, frozen: true, placement: {{type: file, path: base.xyz}}}}
  - {{name: bed, material: grain, radius: 0.5, placement: {{type: file, path: bed.xyz}}}}
{floor}time: {{dt: 1e-4, end: {end}}}
neighbor: {{skin: 0.1}}
output: {{every: {end}}}
""")

with open(work + "/data.chute", "w") as f:
    f.write("chute scene of grains' bench/chute/gen.py\n\n%d atoms\n2 atom types\n\n" % (len(base) + len(bed)))
    f.write("0 %.17g xlo xhi\n0 %.17g ylo yhi\n-1 %.17g zlo zhi\n\nAtoms # sphere\n\n" % (L, L, zmax))
    k = 0
    for p in bed:
        k += 1
        f.write("%d 1 1 1 %.17g %.17g %.17g\n" % ((k,) + p))
    for p in base:
        k += 1
        f.write("%d 2 1 1 %.17g %.17g %.17g\n" % ((k,) + p))

with open(work + "/in.chute", "w") as f:
    f.write("""# grains bench/chute: LAMMPS's chute benchmark on grains' scene
units           lj
atom_style      sphere
boundary        p p fm
newton          off
comm_modify     vel yes
read_data       data.chute
pair_style      gran/hooke/history 200000.0 NULL 50.0 NULL 0.5 0
pair_coeff      * *
neighbor        0.1 bin
neigh_modify    every 1 delay 0
timestep        0.0001
group           bottom type 2
group           active subtract all bottom
neigh_modify    exclude group bottom bottom
fix             1 all gravity 1.0 chute %g
fix             2 bottom freeze
fix             3 active nve/sphere
compute         ke active ke
variable        vx equal vcm(active,x)
thermo_style    custom step atoms c_ke v_vx
thermo_modify   norm no
thermo          %d
run             %d
""" % (angle, steps, steps))
print("N=%d BASE=%d BED=%d L=%g" % (len(base) + len(bed), len(base), len(bed), L))
