#pragma once
// The peak resident memory of this process, per run: Linux keeps the high-water mark
// (VmHWM in /proc/self/status), and writing "5" to /proc/self/clear_refs resets it.

namespace gplan {

// Resets the high-water mark to the current resident size; false where it cannot.
bool reset_peak_memory();
// Peak resident memory since the last reset (or the process start), in MB (2^20
// bytes); NaN where /proc does not say.
double peak_memory_mb();

}  // namespace gplan
