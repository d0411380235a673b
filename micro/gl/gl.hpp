#pragma once
// The one place GL is included from: glad2's generated loader (built by CMake from python3-glad).
#include <glad/gl.h>
