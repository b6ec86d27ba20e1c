#pragma once
// A damaged HDF5 file must never take flag-sim down. libhdf5 trusts the
// metadata it reads (object headers, global heaps, chunk indexes): a few
// flipped bits can send it out of bounds (a SIGSEGV in H5HG_read, reached from
// a variable-length string attribute, or a heap corrupted until free()
// aborts). So the risky reads run in a forked child first:
//  - `info` reads everything it reports in the child and only prints what the
//    child returns (run_isolated): the process that prints never ran a read;
//  - every OutputReader first has a child open the file and make the reads the
//    commands make, in the order they make them, then walk every object and
//    attribute (OutputReader's constructor). The child starts from the same
//    address space as its parent (fork), so a read that crashes the parent
//    crashes the child first, and the file is refused with one error line.
#include <functional>
#include <string>

namespace flagsim::data {

/// Runs `work` in a forked child and returns the string it returned. A
/// UserError or IoError it throws is thrown again here with the same message;
/// a child killed by a signal (or one that could not report) is a UserError
/// naming `path` as damaged. Without fork (no memory for a child), `work` runs here.
std::string run_isolated(const std::string& path, const std::function<std::string()>& work);

/// True inside run_isolated's child: OutputReader does not fork again there.
bool in_isolated_child();

/// Whether OutputReader makes its test read in a child (default true). The
/// output reader's fuzz target turns it off: it wants a crash in our reads to
/// be a crash it sees, and runs the test read's walk in-process instead.
bool isolated_reads();
void set_isolated_reads(bool on);

}  // namespace flagsim::data
