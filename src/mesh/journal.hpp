#pragma once
// Taking changes back, level by level. A local operation is tried and judged afterwards (§4.1: an
// operation is kept only if it improves the energy); a move of the curve stage may need a repair
// made of such operations, judged as a whole (§4.2). So the levels nest: open() starts a level
// inside the current one, rollback() takes back the changes of the innermost level alone, and
// commit() hands them to the enclosing level (which may still take them back) or, at the
// outermost level, forgets them.
//
// The triangle mesh journals its own changes (TriMesh::open_journal); what a stage attaches to
// the mesh — the curve stage's nodes and the data of its edges and triangles — lives in the
// stores below, attached to the mesh's Journal, so that one call takes back the mesh and its
// attributes together and no stage copies anything to undo.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

namespace curvemesh::mesh {

// A store whose changes a Journal can take back: it logs each change while its journal records.
class JournalMember {
 public:
  virtual ~JournalMember() = default;
  virtual std::size_t log_length() const = 0;
  virtual void undo_to(std::size_t length) = 0;  // takes back the changes logged after `length`, newest first
  virtual void forget() = 0;                     // empties the log
};

class Journal {
 public:
  Journal() = default;
  // A copy of a mesh has no attributes attached: its journal starts empty and closed.
  Journal(const Journal&) {}
  Journal& operator=(const Journal&) { return *this; }

  // Members attach and detach while no level is open.
  void attach(JournalMember& member);
  void detach(JournalMember& member);

  void open();
  void commit();
  void rollback();
  bool recording() const { return depth_ > 0; }
  bool has_members() const { return !members_.empty(); }
  int depth() const { return depth_; }

 private:
  std::vector<JournalMember*> members_;
  std::vector<std::size_t> marks_;  // per open level, each member's log length when it opened
  int depth_ = 0;
};

// A vector whose changes its journal can take back. Reading is as from a vector; writing goes
// through set, push_back and resize.
template <class T>
class JournaledVector final : public JournalMember {
 public:
  explicit JournaledVector(Journal& journal) : journal_(journal) { journal_.attach(*this); }
  ~JournaledVector() override { journal_.detach(*this); }
  JournaledVector(const JournaledVector&) = delete;
  JournaledVector& operator=(const JournaledVector&) = delete;

  std::size_t size() const { return values_.size(); }
  const T& operator[](std::size_t i) const { return values_[i]; }
  const std::vector<T>& values() const { return values_; }

  void set(std::size_t i, const T& value) {
    if (journal_.recording()) log_.push_back({i, values_[i]});
    values_[i] = value;
  }
  void push_back(const T& value) {
    if (journal_.recording()) log_.push_back({values_.size(), std::nullopt});
    values_.push_back(value);
  }
  void resize(std::size_t n, const T& fill = T{}) {
    while (values_.size() > n) {
      if (journal_.recording()) log_.push_back({values_.size() - 1, values_.back()});
      values_.pop_back();
    }
    while (values_.size() < n) push_back(fill);
  }
  // Replaces every value; only while nothing records (a stage's set-up and compaction).
  void assign(std::vector<T> values) {
    if (journal_.recording()) throw std::logic_error("JournaledVector::assign while the journal records");
    values_ = std::move(values);
  }

  std::size_t log_length() const override { return log_.size(); }
  void undo_to(std::size_t length) override {
    while (log_.size() > length) {
      Entry& e = log_.back();
      if (!e.old) values_.pop_back();
      else if (e.index == values_.size()) values_.push_back(std::move(*e.old));  // a pop taken back
      else values_[e.index] = std::move(*e.old);
      log_.pop_back();
    }
  }
  void forget() override { log_.clear(); }

 private:
  struct Entry {
    std::size_t index;
    std::optional<T> old;  // what was at `index` (set or popped), or nothing: the entry pushed it
  };
  Journal& journal_;
  std::vector<T> values_;
  std::vector<Entry> log_;
};

// A hash map whose changes its journal can take back.
template <class K, class V>
class JournaledMap final : public JournalMember {
 public:
  explicit JournaledMap(Journal& journal) : journal_(journal) { journal_.attach(*this); }
  ~JournaledMap() override { journal_.detach(*this); }
  JournaledMap(const JournaledMap&) = delete;
  JournaledMap& operator=(const JournaledMap&) = delete;

  bool contains(const K& key) const { return values_.count(key) > 0; }
  const V& at(const K& key) const { return values_.at(key); }
  const V* find(const K& key) const {
    const auto it = values_.find(key);
    return it == values_.end() ? nullptr : &it->second;
  }
  bool empty() const { return values_.empty(); }

  void set(const K& key, const V& value) {
    auto [it, inserted] = values_.try_emplace(key, value);
    if (journal_.recording()) log_.push_back({key, inserted ? std::nullopt : std::optional<V>(it->second)});
    if (!inserted) it->second = value;
  }
  void erase(const K& key) {
    const auto it = values_.find(key);
    if (it == values_.end()) return;
    if (journal_.recording()) log_.push_back({key, std::move(it->second)});
    values_.erase(it);
  }
  // Replaces every entry; only while nothing records.
  void assign(std::unordered_map<K, V> values) {
    if (journal_.recording()) throw std::logic_error("JournaledMap::assign while the journal records");
    values_ = std::move(values);
  }

  std::size_t log_length() const override { return log_.size(); }
  void undo_to(std::size_t length) override {
    while (log_.size() > length) {
      auto& [key, old] = log_.back();
      if (old) values_.insert_or_assign(key, std::move(*old));
      else values_.erase(key);
      log_.pop_back();
    }
  }
  void forget() override { log_.clear(); }

 private:
  Journal& journal_;
  std::unordered_map<K, V> values_;
  std::vector<std::pair<K, std::optional<V>>> log_;
};

}  // namespace curvemesh::mesh
