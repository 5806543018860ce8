// The part of every precompiled header: standard and third-party headers that many translation
// units include and that never change while one works on zraka. No zraka header is here (see
// cmake/ZrakaPch.cmake for why). Only headers whose parse is the cost: including one here must
// not emit code in every translation unit (a namespace-scope object with a constructor would).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <locale>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <bit>

// The SIMD intrinsics of the triangle BVH's traversal (triangle_bvh.hpp): ~0.4 CPU-s of parsing.
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

// The scene file reader's parsers: about a second of parsing for each unit that loads scenes.
#if __has_include(<yaml-cpp/yaml.h>)
#include <yaml-cpp/yaml.h>
#endif
