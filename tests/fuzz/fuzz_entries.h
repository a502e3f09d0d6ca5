/// Fuzz entry points shared by the libFuzzer targets (tests/fuzz/*_fuzz.cpp, `make fuzz`) and
/// the corpus replay test that runs in `make test` (tests/fuzz/corpus_replay_test.cpp).
///
/// Contract: bad input is a UserError, which the entry swallows (Outcome::kRefused). Anything else is
/// a bug and escapes: an InternalError or any other exception (libFuzzer then reports an
/// uncaught exception; the replay test fails), a crash, a sanitizer report, or a violated
/// post-condition (a scene that parses but holds a non-finite number, an image that reads
/// but holds a non-finite pixel or a bad size), which aborts through FuzzFail.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace aalab::fuzz {

/// What an entry made of its input: accepted (parsed or read, post-conditions checked) or
/// refused with a UserError. The corpus replay checks it against the file's name.
enum class Outcome { kAccepted, kRefused };

/// Parses the bytes as a scene file (ParseScene; mesh paths resolve against the scene
/// library folder) and checks that a scene that parses is finite and within its documented
/// ranges.
Outcome CheckSceneBytes(const uint8_t* data, size_t size);

/// Writes bytes 1.. to a temporary file whose extension the first byte picks (.png, .exr,
/// .tif by value % 3; no bytes: refused, there is no file), reads it with ReadImage (pixel
/// limit kFuzzMaxPixels) and checks what a successful read returns.
Outcome CheckImageBytes(const uint8_t* data, size_t size);

/// The libFuzzer entries: CheckSceneBytes / CheckImageBytes, returning 0 (libFuzzer's rule).
int FuzzScene(const uint8_t* data, size_t size);
int FuzzImage(const uint8_t* data, size_t size);

/// ReadImage's pixel limit inside FuzzImage: small, so a header that claims a huge image
/// is refused before the (legitimate, documented) allocation of up to 2^28 pixels.
inline constexpr size_t kFuzzMaxPixels = size_t{1} << 16;

/// Reports a violated post-condition on stderr and aborts (a fuzzer finding).
[[noreturn]] void FuzzFail(const std::string& what);

}  // namespace aalab::fuzz
