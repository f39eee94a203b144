// An OpenGL 3.3 core context with no display at all (EGL on Mesa's surfaceless platform) and a
// multisampled framebuffer to draw into, whose pixels can be read back.
#pragma once

#include <tandem/types.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace tandem::render {

// The bound read framebuffer's (0, 0, width, height) pixels as RGB, top row first.
std::vector<uint8_t> readFramebufferPixels(int width, int height);

class OffscreenTarget {
 public:
  // Makes the context current on this thread. An error says which EGL or GL step failed.
  static Result<std::unique_ptr<OffscreenTarget>> create(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  void bind();  // draw into it (done by create)
  // Resolves the samples and returns width × height RGB pixels, top row first.
  std::vector<uint8_t> readPixels();
  int width() const;
  int height() const;

 private:
  OffscreenTarget();
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace tandem::render
