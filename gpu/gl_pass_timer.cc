#include "gpu/gl_pass_timer.h"

#include <stdexcept>
#include <utility>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"

namespace relief::gpu {

GlPassTimer::GlPassTimer() {
  // GL_ARB_timer_query is core since 3.3, but a GL may still give its counter no bits.
  GLint bits = 0;
  glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
  available_ = bits > 0;
}

GlName& GlPassTimer::query(std::size_t index) {
  while (queries_.size() <= index) {
    GLuint name = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &name);
    queries_.emplace_back(GlName::Kind::kQuery, name, current_egl_context());
  }
  return queries_[index];
}

void GlPassTimer::begin(std::string name) {
  if (!available_) {
    return;
  }
  if (open_) {
    throw std::logic_error("GlPassTimer::begin(" + name + "): the pass " + names_.back() +
                           " has not ended");
  }
  glQueryCounter(query(2 * names_.size()).get(), GL_TIMESTAMP);
  names_.push_back(std::move(name));
  open_ = true;
}

void GlPassTimer::end() {
  if (!available_ || !open_) {
    return;
  }
  glQueryCounter(query(2 * names_.size() - 1).get(), GL_TIMESTAMP);
  open_ = false;
}

std::vector<GlPassTime> GlPassTimer::collect() {
  end();
  std::vector<GlPassTime> passes;
  passes.reserve(names_.size());
  for (std::size_t k = 0; k < names_.size(); ++k) {
    GLuint64 start = 0, stop = 0;
    glGetQueryObjectui64v(queries_[2 * k].get(), GL_QUERY_RESULT, &start);
    glGetQueryObjectui64v(queries_[2 * k + 1].get(), GL_QUERY_RESULT, &stop);
    // Nanoseconds; the counter is monotonic, the guard is for a GL whose counter wraps.
    passes.push_back({std::move(names_[k]), stop >= start ? double(stop - start) * 1e-6 : 0.0});
  }
  names_.clear();
  return passes;
}

void GlPassTimer::clear() {
  names_.clear();
  open_ = false;
}

}  // namespace relief::gpu
