// EGL surfaceless context and framebuffers for rendering with no display.
#include "render/offscreen.h"

#include "render/gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

namespace tandem::render {

struct OffscreenTarget::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  int width = 0, height = 0;
  GLuint multisampled = 0, colour = 0, depth = 0;  // framebuffer with 4 samples, colour and depth
  GLuint resolved = 0, resolvedColour = 0;         // one sample, for reading

  ~Impl() {
    if (context != EGL_NO_CONTEXT) {
      glDeleteFramebuffers(1, &multisampled);
      glDeleteFramebuffers(1, &resolved);
      GLuint buffers[] = {colour, depth, resolvedColour};
      glDeleteRenderbuffers(3, buffers);
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    if (display != EGL_NO_DISPLAY) eglTerminate(display);
  }
};

std::vector<uint8_t> readFramebufferPixels(int width, int height) {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<uint8_t> upsideDown(static_cast<size_t>(width) * height * 3);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, upsideDown.data());
  std::vector<uint8_t> pixels(upsideDown.size());  // GL's first row is the bottom one
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(upsideDown.begin() + static_cast<long>((height - 1 - y) * row), row,
                pixels.begin() + static_cast<long>(y * row));
  return pixels;
}

OffscreenTarget::OffscreenTarget() : m_impl(std::make_unique<Impl>()) {}
OffscreenTarget::~OffscreenTarget() = default;

namespace {
Error eglError(const std::string& what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", eglGetError());
  return Error{"offscreen rendering: " + what + " failed (EGL error " + code +
               "); it needs Mesa's EGL (Debian: libegl-mesa0, libgl1-mesa-dri)"};
}
}  // namespace

Result<std::unique_ptr<OffscreenTarget>> OffscreenTarget::create(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    return Error{"offscreen rendering: size must be 1 to 16384 pixels a side, got " + std::to_string(width) + "x" +
                 std::to_string(height)};
  std::unique_ptr<OffscreenTarget> target(new OffscreenTarget());
  Impl& t = *target->m_impl;
  t.width = width;
  t.height = height;
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) return eglError("finding eglGetPlatformDisplayEXT");
  t.display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (t.display == EGL_NO_DISPLAY || !eglInitialize(t.display, &major, &minor))
    return eglError("opening the surfaceless display");
  if (!eglBindAPI(EGL_OPENGL_API)) return eglError("binding OpenGL");
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  t.context = eglCreateContext(t.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, contextAttributes);
  if (t.context == EGL_NO_CONTEXT) return eglError("creating an OpenGL 3.3 core context");
  if (!eglMakeCurrent(t.display, EGL_NO_SURFACE, EGL_NO_SURFACE, t.context)) return eglError("making it current");

  auto makeFramebuffer = [&](GLuint& framebuffer, GLuint& colourBuffer, GLuint* depthBuffer, int samples) {
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glGenRenderbuffers(1, &colourBuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, colourBuffer);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colourBuffer);
    if (depthBuffer) {
      glGenRenderbuffers(1, depthBuffer);
      glBindRenderbuffer(GL_RENDERBUFFER, *depthBuffer);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, *depthBuffer);
    }
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  };
  if (!makeFramebuffer(t.resolved, t.resolvedColour, nullptr, 0) ||
      !makeFramebuffer(t.multisampled, t.colour, &t.depth, 4))
    return Error{"offscreen rendering: the framebuffer is incomplete"};
  return target;
}

void OffscreenTarget::bind() { glBindFramebuffer(GL_FRAMEBUFFER, m_impl->multisampled); }

std::vector<uint8_t> OffscreenTarget::readPixels() {
  const Impl& t = *m_impl;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.multisampled);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.resolved);
  glBlitFramebuffer(0, 0, t.width, t.height, 0, 0, t.width, t.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.resolved);
  std::vector<uint8_t> pixels = readFramebufferPixels(t.width, t.height);
  glBindFramebuffer(GL_FRAMEBUFFER, t.multisampled);
  return pixels;
}

int OffscreenTarget::width() const { return m_impl->width; }
int OffscreenTarget::height() const { return m_impl->height; }

}  // namespace tandem::render
