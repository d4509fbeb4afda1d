#pragma once
// What a number field shows for a value. A pose re-expressed for a new pivot or mirrored for a
// twin leaves components like -1e-17, which "%.4f" prints as "-0.0000": a sign on nothing.

namespace primo::editor {

// `value`, or +0 where it prints as zero with `decimals` places (|value| below half a unit of
// the last place).
double shown_value(double value, int decimals);

}  // namespace primo::editor
