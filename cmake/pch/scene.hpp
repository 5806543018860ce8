// The precompiled header of the programs that render scenes (a chapter or benchmark whose sources
// include one of the headers below, see zraka_pch_kind in cmake/ZrakaPch.cmake): the common part
// plus zraka's scene-level headers, whose parsing was most of such a unit's front end.
// Measured (tools/build_times.sh, touch main.cpp): 2.3-pathtrace 2.39 -> 1.77 s, 6.4-metropolis
// 2.76 -> 2.09 s. The earlier programs (1.0-1.6, 3.1, ...) keep programs.hpp: they include few
// of these headers, and loading this larger PCH would cost them more than it saves.
#pragma once
#include "common.hpp"

#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/app/reference.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>
