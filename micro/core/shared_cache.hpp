#pragma once
// What the cases of one run can share instead of each building its own copy: a scene's meshes for a view
// (the engine grid's 12.76 M triangles take ~13 s to generate and upload on llvmpipe, and a paired
// baseline is prepared once per interleaved group). Owned by the runner, so nothing outlives the GL
// context; reached through CaseContext::shared(). Entries are keyed by text (the builder names everything
// the value depends on) and by type; of each type the `capacity` most recently used stay (a type of small
// values may keep more: get()'s `keep`), and a case keeps what it got alive after that (shared_ptr), so
// memory is bounded by the live cases plus the capacity per type.
#include <cstddef>
#include <functional>
#include <list>
#include <memory>
#include <string>
#include <typeinfo>

namespace oitbench {

class SharedCache {
 public:
  explicit SharedCache(size_t capacity = 2) : capacity_(capacity) {}
  SharedCache(const SharedCache&) = delete;
  SharedCache& operator=(const SharedCache&) = delete;

  // The value stored under `key`, or make()'s, stored (a make() that throws stores nothing). `keep`: the
  // most entries of type T kept (0: the cache's capacity), for small values many cases share (a pool's
  // size) beside big ones (a scene's meshes); each type's entries are evicted only by its own kind.
  template <class T>
  std::shared_ptr<const T> get(const std::string& key, const std::function<std::shared_ptr<const T>()>& make,
                               size_t keep = 0) {
    const std::string type = std::string(typeid(T).name()) + '\n';
    const std::string full = type + key;
    for (auto it = entries_.begin(); it != entries_.end(); ++it)
      if (it->key == full) {
        entries_.splice(entries_.begin(), entries_, it);
        ++hits_;
        return std::static_pointer_cast<const T>(entries_.front().value);
      }
    std::shared_ptr<const T> made = make();
    ++misses_;
    if (capacity_ == 0) return made;
    entries_.push_front({full, made});
    size_t of_type = 0;
    for (auto it = entries_.begin(); it != entries_.end();)
      if (it->key.compare(0, type.size(), type) == 0 && ++of_type > (keep ? keep : capacity_))
        it = entries_.erase(it);
      else
        ++it;
    return made;
  }
  unsigned hits() const { return hits_; }
  unsigned misses() const { return misses_; }

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const void> value;
  };
  size_t capacity_;
  std::list<Entry> entries_;  // most recently used first
  unsigned hits_ = 0, misses_ = 0;
};

}  // namespace oitbench
