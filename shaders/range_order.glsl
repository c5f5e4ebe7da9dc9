// The automatic ranges' order of floats (view_range.comp, view_decode.comp); its inverse on the CPU
// is views/ui/view_map.h floatFromOrdered.

// Monotonic map of floats to uints (negative floats below positive ones), so atomicMin/Max work.
uint orderedFromFloat(float f) {
  uint b = floatBitsToUint(f);
  return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}
