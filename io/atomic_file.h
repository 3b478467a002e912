#pragma once

#include <filesystem>
#include <functional>
#include <vector>

namespace clipblur {

// Several files replaced as one: write() fills a temporary beside each target, and commit() renames
// them over their targets, in the order written, only once every write has succeeded. A failed write
// throws and a group destroyed uncommitted removes its temporaries, so the previous targets are all
// untouched. commit() first refuses targets that became folders, the one rename failure a pre-render
// check of the output paths cannot rule out for good; a rename failing after that (the disk itself)
// leaves the files already renamed in place. Errors are clipblur::Error (ExitCode::Output).
class AtomicFileGroup {
public:
    using Writer = std::function<void(const std::filesystem::path& temporary)>;

    AtomicFileGroup() = default;
    AtomicFileGroup(const AtomicFileGroup&) = delete;
    AtomicFileGroup& operator=(const AtomicFileGroup&) = delete;
    ~AtomicFileGroup();

    void write(const std::filesystem::path& target, const Writer& write);
    void commit();

private:
    struct Pending {
        std::filesystem::path target;
        std::filesystem::path temporary;
    };
    std::vector<Pending> pending_;
};

// One file written all or nothing: a group of one, committed.
void writeAtomically(const std::filesystem::path& target, const AtomicFileGroup::Writer& write);

}  // namespace clipblur
