#pragma once
// The version and the commit this build was made from (`dtlab --version`, dtlab.__version__).

namespace dtlab {

const char* version();       // the project's version, e.g. "0.1.0"
const char* build_commit();  // the full commit hash, "+uncommitted" when the tree had changes

}  // namespace dtlab
