#pragma once
// Quality metrics as `primo metrics` and `primo bench quality` report them: the same JSON keys
// and the same number formats in both.

#include <nlohmann/json.hpp>
#include <string>

#include "mesh_quality.h"

namespace primo::quality {

// Every field of the metrics; volume_change_percent is null when the rest volume is zero.
nlohmann::json quality_json(const QualityMetrics& metrics);

// "+12.3" (one decimal, signed), or "-" when the rest volume is zero.
std::string format_volume_change(const QualityMetrics& metrics);

}  // namespace primo::quality
