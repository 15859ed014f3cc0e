// SPDX-License-Identifier: MIT
// The translation unit that builds the tests' precompiled header (tests/CMakeLists.txt,
// smi_test_pch): Catch2 and Eigen's dense module, which nearly every test program includes.
