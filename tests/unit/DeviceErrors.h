// The fixtures of the device-error suites, shared by the *ErrorTests.cpp files (one topic each).
#pragma once
#include <array>
#include <atomic>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <thread>
#include <gtest/gtest.h>

#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/ShaderReflection.h"
#include "fe/gdi/ShaderRegistry.h"
#include "fe/gdi/Validation.h"

// Mistakes made through the device on every backend: the same gdi::Error before any native call.
class DeviceErrors : public fe::testing::BackendTest {};
// Damaged SPIR-V is refused by createShader with an Error naming the shader, on every backend;
// before SPIR-V was validated, SPIRV-Cross's reflection crashed on some such modules (found by
// the capture-file fuzzer).
class DamagedSpirv : public fe::testing::BackendTest {};
