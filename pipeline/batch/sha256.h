#pragma once
// SHA-256 (FIPS 180-4): the content keys of batch variants and the digests
// of their output files. No crypto library is among the project's
// dependencies; this one is checked against the FIPS 180-2 test vectors.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace fabmesh {

/// Whether this processor has the x86 SHA extensions (SHA-NI) that
/// Sha256 uses when it may.
bool sha256_hardware();

/// An incremental SHA-256: update() any number of times, then digest().
/// The blocks are compressed with the x86 SHA extensions where the
/// processor has them (about eight times faster), else portably; the
/// digests are the same.
class Sha256 {
 public:
  enum class Engine {
    Fastest,   ///< the SHA extensions when the processor has them
    Portable,  ///< the portable code always (the tests compare the two)
  };
  explicit Sha256(Engine engine = Engine::Fastest);
  /// Adds `bytes` to the message.
  Sha256& update(std::string_view bytes);
  /// The 32-byte digest of everything added; the object must not be updated afterwards.
  std::array<std::uint8_t, 32> digest();
  /// digest() as 64 lowercase hexadecimal digits.
  std::string hex_digest();

 private:
  void compress(const std::uint8_t* blocks, std::size_t count);

  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;  ///< message length in bytes
  bool hardware_ = false;     ///< compress with the SHA extensions
};

/// The SHA-256 of `bytes` as 64 lowercase hexadecimal digits.
std::string sha256_hex(std::string_view bytes);

}  // namespace fabmesh
