#include "shown_value.h"

#include <cmath>

namespace primo::editor {

double shown_value(double value, int decimals) {
  return std::abs(value) < 0.5 * std::pow(10.0, -decimals) ? 0.0 : value;
}

}  // namespace primo::editor
