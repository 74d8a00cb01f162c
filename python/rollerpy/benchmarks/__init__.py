"""The runners of the C++ benchmark programs in benchmarks/ (docs/benchmarks.md), each a command."""
