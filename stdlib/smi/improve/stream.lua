--- smi.improve.stream(seed, label) -> seed: the integer seed of the study's random stream named
-- `label` (smi.rng's named streams), for the kernels that take an integer seed. Each random step
-- of a study draws from its own stream of the study's seed, so a new step changes no other
-- step's numbers, and no two steps share a sequence by a coincidence of hand-picked offsets.
return function(seed, label)
  return math.tointeger(smi.rng(seed, label):integers(1, 0, 2147483646)[1])
end
