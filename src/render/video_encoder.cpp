#include "render/video_encoder.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <unistd.h>

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "common/stop.h"

namespace aerobox {

struct VideoEncoder::Impl {
  std::string path;
  std::string partial;
  int width = 0;
  int height = 0;
  int fps = 0;
  size_t capacity = 8;

  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scale = nullptr;
  bool header_written = false;
  bool finished = false;

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Image> queue;
  bool closing = false;
  std::string error;  // the worker's failure, if any
  int written = 0;
  std::thread worker;

  void Check(int code, const char* what) {
    if (code < 0) {
      char text[AV_ERROR_MAX_STRING_SIZE] = {0};
      av_strerror(code, text, sizeof(text));
      throw std::runtime_error(std::string("video: ") + what + ": " + text);
    }
  }

  // Sends one frame (or nullptr to flush) and writes every packet that comes out.
  void Encode(AVFrame* input) {
    Check(avcodec_send_frame(codec, input), "encoding a frame");
    while (true) {
      if (input == nullptr) ThrowIfStopRequested("encoding the video (its last frames)");
      const int code = avcodec_receive_packet(codec, packet);
      if (code == AVERROR(EAGAIN) || code == AVERROR_EOF) return;
      Check(code, "receiving a packet");
      // the duration must be set before the timestamps are rescaled to the stream's base
      packet->duration = 1;
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      Check(av_interleaved_write_frame(format, packet), "writing a packet");
    }
  }

  void Convert(const Image& image, int64_t index) {
    Check(av_frame_make_writable(frame), "preparing a frame");
    const uint8_t* source[1] = {image.rgb.data()};
    const int stride[1] = {3 * width};
    sws_scale(scale, source, stride, 0, height, frame->data, frame->linesize);
    frame->pts = index;
  }

  void Run() {
    while (true) {
      Image image;
      {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [this] { return !queue.empty() || closing; });
        if (queue.empty()) return;
        if (StopRequested()) {
          // Ctrl-C: the frames still queued are dropped; AddFrame() and Finish() throw
          // Interrupted
          closing = true;
          lock.unlock();
          changed.notify_all();
          return;
        }
        image = std::move(queue.front());
        queue.pop_front();
      }
      changed.notify_all();
      try {
        Convert(image, written);
        Encode(frame);
        std::lock_guard<std::mutex> lock(mutex);
        ++written;
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex);
        error = e.what();
        queue.clear();
        closing = true;
        changed.notify_all();
        return;
      }
    }
  }

  void StopWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      closing = true;
    }
    changed.notify_all();
    if (worker.joinable()) worker.join();
  }

  void Release() {
    // each pointer is cleared as it is freed: Release() runs again from the destructor when
    // Finish() failed after releasing (a rename that did not succeed)
    sws_freeContext(scale);
    scale = nullptr;
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (format != nullptr) {
      if (format->pb != nullptr) avio_closep(&format->pb);
      avformat_free_context(format);
      format = nullptr;
    }
  }
};

VideoEncoder::VideoEncoder(const std::string& path, int width, int height, int fps,
                           int queue_capacity)
    : impl_(std::make_unique<Impl>()) {
  Impl& v = *impl_;
  if (width % 2 != 0 || height % 2 != 0 || width <= 0 || height <= 0) {
    throw std::runtime_error("video: width and height must be even and positive for yuv420p");
  }
  if (fps <= 0) throw std::runtime_error("video: fps must be positive");
  av_log_set_level(AV_LOG_ERROR);
  v.path = path;
  v.partial = TemporaryPath(path);
  v.width = width;
  v.height = height;
  v.fps = fps;
  v.capacity = static_cast<size_t>(std::max(1, queue_capacity));
  try {
    v.Check(avformat_alloc_output_context2(&v.format, nullptr, "mp4", v.partial.c_str()),
            "creating the MP4 container");
    const AVCodec* h264 = avcodec_find_encoder_by_name("libx264");
    if (h264 == nullptr) h264 = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (h264 == nullptr) throw std::runtime_error("video: no H.264 encoder in this libavcodec");
    v.stream = avformat_new_stream(v.format, nullptr);
    v.codec = avcodec_alloc_context3(h264);
    if (v.stream == nullptr || v.codec == nullptr) throw std::runtime_error("video: out of memory");
    v.codec->width = width;
    v.codec->height = height;
    v.codec->pix_fmt = AV_PIX_FMT_YUV420P;
    v.codec->time_base = AVRational{1, fps};
    v.codec->framerate = AVRational{fps, 1};
    v.codec->gop_size = 2 * fps;
    if (v.format->oformat->flags & AVFMT_GLOBALHEADER)
      v.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    av_opt_set(v.codec->priv_data, "preset", "veryfast", 0);
    av_opt_set(v.codec->priv_data, "crf", "23", 0);
    v.Check(avcodec_open2(v.codec, h264, nullptr), "opening the H.264 encoder");
    v.Check(avcodec_parameters_from_context(v.stream->codecpar, v.codec), "describing the stream");
    v.stream->time_base = v.codec->time_base;
    v.Check(avio_open(&v.format->pb, v.partial.c_str(), AVIO_FLAG_WRITE), "opening the file");
    AVDictionary* options = nullptr;
    av_dict_set(&options, "movflags", "+faststart", 0);
    const int header = avformat_write_header(v.format, &options);
    av_dict_free(&options);
    v.Check(header, "writing the header");
    v.header_written = true;
    v.frame = av_frame_alloc();
    v.packet = av_packet_alloc();
    if (v.frame == nullptr || v.packet == nullptr) throw std::runtime_error("video: out of memory");
    v.frame->format = AV_PIX_FMT_YUV420P;
    v.frame->width = width;
    v.frame->height = height;
    v.Check(av_frame_get_buffer(v.frame, 0), "allocating a frame");
    v.scale = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P,
                             SWS_BILINEAR, nullptr, nullptr, nullptr);
    if (v.scale == nullptr) throw std::runtime_error("video: no RGB to YUV converter");
  } catch (...) {
    v.Release();
    std::remove(v.partial.c_str());
    throw;
  }
  v.worker = std::thread([this] { impl_->Run(); });
}

VideoEncoder::~VideoEncoder() {
  Impl& v = *impl_;
  v.StopWorker();
  if (!v.finished) {
    v.Release();
    std::remove(v.partial.c_str());
  }
}

void VideoEncoder::AddFrame(Image frame) {
  Impl& v = *impl_;
  if (frame.width != v.width || frame.height != v.height) {
    throw std::runtime_error("video: frame size differs from the video's");
  }
  std::unique_lock<std::mutex> lock(v.mutex);
  v.changed.wait(lock,
                 [&v] { return v.queue.size() < v.capacity || !v.error.empty() || v.closing; });
  if (!v.error.empty()) throw std::runtime_error(v.error);
  if (v.closing) ThrowIfStopRequested("encoding the video");
  v.queue.push_back(std::move(frame));
  lock.unlock();
  v.changed.notify_all();
}

void VideoEncoder::Finish() {
  Impl& v = *impl_;
  v.StopWorker();  // drains the queue first: the worker leaves only when it is empty
  if (!v.error.empty()) throw std::runtime_error(v.error);
  ThrowIfStopRequested("encoding the video");
  v.Encode(nullptr);  // flush
  v.Check(av_write_trailer(v.format), "writing the trailer");
  v.Release();
  if (std::rename(v.partial.c_str(), v.path.c_str()) != 0) {
    std::remove(v.partial.c_str());
    throw std::runtime_error("video: cannot move " + v.partial + " into place");
  }
  v.finished = true;
}

std::string VideoEncoder::TemporaryPath(const std::string& path) {
  return path + "." + std::to_string(getpid()) + ".partial";
}

int VideoEncoder::frames_written() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->written;
}

}  // namespace aerobox
