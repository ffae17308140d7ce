// The one Catch2 main, compiled once per build and linked into every test
// binary (the Catch2 2 header is slow to compile).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
