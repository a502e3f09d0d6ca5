// libFuzzer target: image files (ReadImage on PNG/EXR/TIFF by the first byte). Built and run by
// `make fuzz` (scripts/fuzz.sh).
#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return aalab::fuzz::FuzzImage(data, size); }
