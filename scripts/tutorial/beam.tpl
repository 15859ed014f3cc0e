# smi-beam-solver input deck, written by smi-lua from beam.tpl for one point
E   = {{E}}     # Young's modulus, MPa
h   = {{h}}     # thickness, mm
b   = {{b}}     # width, mm
L   = {{L}}     # free length, mm
rho = 7.85e-9   # density, t/mm^3 (steel)
