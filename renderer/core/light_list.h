// Scene::lights: the point lights, with a generation number that every non-const access changes,
// so the renderer can tell in O(1) whether the lights may differ from what it uploaded (light
// setup on the GPU, renderer/gpu/gpu_lights.cpp) instead of comparing every light each frame.
#pragma once
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

#include "renderer/core/lights.h"

namespace gb {

// A vector of lights whose non-const members (element access, iterators, data(), every edit,
// assignment) each draw a new generation from one process-wide counter before returning, so a
// copy, a moved-from list and a list of another scene never share one. Const access leaves it.
// A reference or iterator obtained through non-const access is for edits before the next frame
// is rendered: an edit through one kept across a frame would not be seen (with validation on, the
// renderer compares the lights anyway and stops on such an edit: gpu_lights.cpp).
class LightList {
 public:
  using Vector = std::vector<PointLightDesc>;
  using value_type = PointLightDesc;
  using size_type = std::size_t;
  using iterator = Vector::iterator;
  using const_iterator = Vector::const_iterator;
  using reference = PointLightDesc&;
  using const_reference = const PointLightDesc&;

  LightList() : gen_(nextGeneration()) {}
  LightList(Vector v) : v_(std::move(v)), gen_(nextGeneration()) {}  // NOLINT: a vector converts
  LightList(std::initializer_list<PointLightDesc> l) : v_(l), gen_(nextGeneration()) {}
  explicit LightList(size_type n, const PointLightDesc& value = {}) : v_(n, value), gen_(nextGeneration()) {}
  LightList(const LightList& o) : v_(o.v_), gen_(nextGeneration()) {}
  LightList(LightList&& o) noexcept : v_(std::move(o.v_)), gen_(nextGeneration()) { o.touch(); }
  LightList& operator=(const LightList& o) { return v_ = o.v_, touched(); }
  LightList& operator=(LightList&& o) noexcept { return v_ = std::move(o.v_), o.touch(), touched(); }
  LightList& operator=(Vector v) { return v_ = std::move(v), touched(); }
  LightList& operator=(std::initializer_list<PointLightDesc> l) { return v_ = l, touched(); }

  // ---- const access: the generation stays ----
  uint64_t generation() const { return gen_; }
  size_type size() const { return v_.size(); }
  bool empty() const { return v_.empty(); }
  const PointLightDesc& operator[](size_type i) const { return v_[i]; }
  const PointLightDesc& at(size_type i) const { return v_.at(i); }
  const PointLightDesc& front() const { return v_.front(); }
  const PointLightDesc& back() const { return v_.back(); }
  const_iterator begin() const { return v_.begin(); }
  const_iterator end() const { return v_.end(); }
  const_iterator cbegin() const { return v_.cbegin(); }
  const_iterator cend() const { return v_.cend(); }
  const PointLightDesc* data() const { return v_.data(); }
  const Vector& vector() const { return v_; }
  operator const Vector&() const { return v_; }  // NOLINT: reads as the vector it wraps

  // ---- non-const access: a new generation, then the access ----
  PointLightDesc& operator[](size_type i) { return touch(), v_[i]; }
  PointLightDesc& at(size_type i) { return touch(), v_.at(i); }
  PointLightDesc& front() { return touch(), v_.front(); }
  PointLightDesc& back() { return touch(), v_.back(); }
  iterator begin() { return touch(), v_.begin(); }
  iterator end() { return touch(), v_.end(); }
  PointLightDesc* data() { return touch(), v_.data(); }
  void push_back(const PointLightDesc& l) { touch(), v_.push_back(l); }
  template <class... Args>
  PointLightDesc& emplace_back(Args&&... args) {
    return touch(), v_.emplace_back(std::forward<Args>(args)...);
  }
  void pop_back() { touch(), v_.pop_back(); }
  void assign(size_type n, const PointLightDesc& l) { touch(), v_.assign(n, l); }
  template <class It>
  void assign(It first, It last) { touch(), v_.assign(first, last); }
  void assign(std::initializer_list<PointLightDesc> l) { touch(), v_.assign(l); }
  void resize(size_type n) { touch(), v_.resize(n); }
  void resize(size_type n, const PointLightDesc& l) { touch(), v_.resize(n, l); }
  void clear() { touch(), v_.clear(); }
  void reserve(size_type n) { touch(), v_.reserve(n); }
  iterator erase(const_iterator pos) { return touch(), v_.erase(pos); }
  iterator erase(const_iterator first, const_iterator last) { return touch(), v_.erase(first, last); }
  iterator insert(const_iterator pos, const PointLightDesc& l) { return touch(), v_.insert(pos, l); }
  template <class It>
  iterator insert(const_iterator pos, It first, It last) {
    return touch(), v_.insert(pos, first, last);
  }
  void swap(LightList& o) noexcept { v_.swap(o.v_), touch(), o.touch(); }

 private:
  static uint64_t nextGeneration();  // the process-wide counter (light_list.cpp), atomic
  void touch() { gen_ = nextGeneration(); }
  LightList& touched() { return touch(), *this; }

  Vector v_;
  uint64_t gen_;
};

}  // namespace gb
