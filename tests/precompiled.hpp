// The headers most test files include, compiled once per build folder and handed to every test
// file as a precompiled header (tests/CMakeLists.txt, target_precompile_headers). Parsing them was
// a third to a half of compiling a short test file, in each of CI's builds that compile the tests.
// Only headers most test files include anyway belong here: a test file still includes what it
// uses, so it compiles without this header too (MECHGRAPH_TEST_PCH=OFF).
#pragma once

#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>
