// An OSMesa (CPU) OpenGL context that owns its colour buffer: created current, destroyed with
// the object. MuJoCo's renderer draws into its own off-screen framebuffer inside it.
#pragma once

#include <memory>

namespace aerobox {

// Mesa writes compiled shaders to a disk cache (~/.cache) from a thread of its own, which holds
// up the end of the process: on a loaded machine, a Ctrl-C while a context was being made
// took 0.6-0.9 s to end the process, that thread still running. Turns the cache off, unless
// the user chose otherwise (MESA_SHADER_CACHE_DISABLE set); making a context is as fast without
// it (mjr_makeContext about 0.3 s either way). Call at start-up, before any thread is started.
void DisableShaderDiskCache();

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
