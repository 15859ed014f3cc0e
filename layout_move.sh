#!/usr/bin/env bash
# One-off layout move (deleted after use): infrastructure out of kernels/, file names matching headers.
set -euo pipefail
cd /work/main
mkdir -p host/platform tests/platform
git mv host/kernels/core host/platform/core
git mv host/kernels/eval host/platform/eval
git mv tests/kernels/core tests/platform/core
git mv tests/kernels/eval tests/platform/eval
# Implementation files named after the header they implement (<header>.cpp or <header>_<part>.cpp).
mv_impl() { git mv "$1" "$2"; }
S=host/kernels/surrogate
mv_impl $S/fit.cpp $S/kriging_fit.cpp
mv_impl $S/loo.cpp $S/kriging_loo.cpp
mv_impl $S/predict.cpp $S/kriging_predict.cpp
mv_impl $S/predict_gradient.cpp $S/kriging_predict_gradient.cpp
mv_impl $S/model_io.cpp $S/kriging_model_io.cpp
mv_impl $S/lhs.cpp $S/doe_lhs.cpp
mv_impl $S/sobol.cpp $S/doe_sobol.cpp
mv_impl $S/sobol_indices.cpp $S/screen_sobol_indices.cpp
mv_impl host/kernels/improve/objective_gradient.cpp host/kernels/improve/statistical_objective_gradient.cpp
mv_impl host/sandbox/files.cpp host/sandbox/sandbox_files.cpp
mv_impl host/sandbox/environment.cpp host/sandbox/sandbox_environment.cpp
mv_impl host/luax/vec_mat.cpp host/luax/luax_vec_mat.cpp
mv_impl host/cli/libs_install.cpp host/cli/commands_libs_install.cpp
mv_impl host/cli/libs_pack.cpp host/cli/commands_libs_pack.cpp
# Paths in every tracked text file (includes, comments, docs, scripts, CMake).
files=$(git ls-files | grep -vE '\.(png|svg|gz|tar|bin|xlsx)$' | grep -v '^bench/fuzz_corpus/')
sed -i -E \
  -e 's#kernels/core\b#platform/core#g' -e 's#kernels/eval\b#platform/eval#g' \
  -e 's#surrogate/fit\.cpp#surrogate/kriging_fit.cpp#g' -e 's#surrogate/loo\.cpp#surrogate/kriging_loo.cpp#g' \
  -e 's#surrogate/predict\.cpp#surrogate/kriging_predict.cpp#g' -e 's#surrogate/predict_gradient\.cpp#surrogate/kriging_predict_gradient.cpp#g' \
  -e 's#surrogate/model_io\.cpp#surrogate/kriging_model_io.cpp#g' -e 's#surrogate/lhs\.cpp#surrogate/doe_lhs.cpp#g' \
  -e 's#surrogate/sobol\.cpp#surrogate/doe_sobol.cpp#g' -e 's#surrogate/sobol_indices\.cpp#surrogate/screen_sobol_indices.cpp#g' \
  -e 's#improve/objective_gradient\.cpp#improve/statistical_objective_gradient.cpp#g' \
  -e 's#sandbox/files\.cpp#sandbox/sandbox_files.cpp#g' -e 's#sandbox/environment\.cpp#sandbox/sandbox_environment.cpp#g' \
  -e 's#luax/vec_mat\.cpp#luax/luax_vec_mat.cpp#g' -e 's#cli/libs_install\.cpp#cli/commands_libs_install.cpp#g' \
  -e 's#cli/libs_pack\.cpp#cli/commands_libs_pack.cpp#g' \
  $files
# Runtime lives in app's namespace.
sed -i -E 's/namespace smi::vm \{/namespace smi::app {/; s/\}  \/\/ namespace smi::vm/}  \/\/ namespace smi::app/' host/app/*.cpp host/app/*.hpp
sed -i -E 's/\bvm::(Runtime|Config|default_out_dir)\b/app::\1/g' $(git ls-files 'host/cli/*' 'host/repl/*' 'tests/*.cpp' 'bench/*.cpp')
