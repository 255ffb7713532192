// The headers nearly every mrloc translation unit reads, precompiled once per target
// (MRLOC_PCH, on by default): MRPT's and Eigen's headers are about 6 s of an 8 s compile, and
// CI builds the project twice on two cores. Only third-party and standard headers belong here:
// each source still includes what it uses, so a build with -DMRLOC_PCH=OFF is the check.
#pragma once
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <nlohmann/json.hpp>
