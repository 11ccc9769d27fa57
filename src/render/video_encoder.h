// H.264 MP4 video (yuv420p, faststart) with libavcodec/libavformat, encoded on a worker thread
// fed through a bounded queue, so rendering and encoding overlap. The file is written under a
// temporary name and renamed when finished: it is complete or absent, never corrupt.
#pragma once

#include <memory>
#include <string>

#include "render/image.h"

namespace aerobox {

class VideoEncoder {
 public:
  // Throws std::runtime_error when the encoder or the file cannot be set up; width and height
  // must be even (yuv420p).
  VideoEncoder(const std::string& path, int width, int height, int fps, int queue_capacity = 8);
  // Without Finish(), stops the worker and removes the temporary file.
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // Queues a frame (blocks while the queue is full). Throws std::runtime_error when the worker
  // failed (the reason is in the message) or the frame has the wrong size.
  void AddFrame(Image frame);

  // Drains the queue, flushes the encoder, writes the trailer and renames the file into place.
  void Finish();

  int frames_written() const;

  // The temporary file a video for `path` is written to: "<path>.<process id>.partial", so
  // that two processes never share one.
  static std::string TemporaryPath(const std::string& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aerobox
