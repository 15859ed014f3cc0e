-- SPDX-License-Identifier: MIT
-- A first study in ten lines: characterize nine measurements (placeholder until the
-- steering-column study lands).
local x = smi.vec{30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}
print(("n = %d, mean = %.4f Hz, sd = %.4f Hz"):format(#x, x:mean(), x:std()))
print(("quartiles: %.3f %.3f %.3f"):format(x:quantile(0.25), x:median(), x:quantile(0.75)))
