#include "render/offscreen_context.h"

#include <GL/osmesa.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace aerobox {

void DisableShaderDiskCache() { setenv("MESA_SHADER_CACHE_DISABLE", "true", /*overwrite=*/0); }

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;
  int width = 0;
  int height = 0;
};

OffscreenContext::OffscreenContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  // RGBA, 24-bit depth, 8-bit stencil (MuJoCo uses both)
  impl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (impl_->context == nullptr) throw std::runtime_error("OSMesa could not create a context");
  impl_->width = width;
  impl_->height = height;
  impl_->buffer.resize(static_cast<size_t>(width) * height * 4);
  MakeCurrent();
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context != nullptr) OSMesaDestroyContext(impl_->context);
}

void OffscreenContext::MakeCurrent() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, impl_->width,
                         impl_->height)) {
    throw std::runtime_error("OSMesa could not make its context current (" +
                             std::to_string(impl_->width) + "x" + std::to_string(impl_->height) +
                             ")");
  }
}

void OffscreenContext::ReleaseCurrent() { OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0); }

}  // namespace aerobox
