#include "mesh/journal.hpp"

#include <algorithm>

namespace curvemesh::mesh {

void Journal::attach(JournalMember& member) {
  if (recording()) throw std::logic_error("Journal::attach while a level is open");
  members_.push_back(&member);
}

void Journal::detach(JournalMember& member) {
  // A member leaving with levels open (a stage unwinding from an exception) takes its log along;
  // the other members' marks keep their places.
  const auto it = std::find(members_.begin(), members_.end(), &member);
  if (it == members_.end()) return;
  const std::size_t k = static_cast<std::size_t>(it - members_.begin()), n = members_.size();
  for (std::size_t level = depth_; level-- > 0;) marks_.erase(marks_.begin() + static_cast<std::ptrdiff_t>(level * n + k));
  members_.erase(it);
}

void Journal::open() {
  for (const JournalMember* m : members_) marks_.push_back(m->log_length());
  ++depth_;
}

void Journal::commit() {
  if (depth_ == 0) throw std::logic_error("Journal::commit with no open level");
  marks_.resize(marks_.size() - members_.size());
  if (--depth_ == 0)
    for (JournalMember* m : members_) m->forget();
}

void Journal::rollback() {
  if (depth_ == 0) throw std::logic_error("Journal::rollback with no open level");
  const std::size_t first = marks_.size() - members_.size();
  for (std::size_t k = 0; k < members_.size(); ++k) members_[k]->undo_to(marks_[first + k]);
  marks_.resize(first);
  --depth_;
}

}  // namespace curvemesh::mesh
