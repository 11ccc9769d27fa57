// An OSMesa (CPU) OpenGL context that owns its colour buffer: created current, destroyed with
// the object. MuJoCo's renderer draws into its own off-screen framebuffer inside it.
#pragma once

#include <memory>

namespace aerobox {

class OffscreenContext {
 public:
  // Throws std::runtime_error when OSMesa cannot create or activate a context.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  // Makes this context current on the calling thread.
  void MakeCurrent();
  // Unbinds the calling thread's current context, so that another thread may make this one
  // current (a context is current in at most one thread).
  static void ReleaseCurrent();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aerobox
