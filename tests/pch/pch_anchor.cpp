// The precompiled headers of the tests (tests/CMakeLists.txt) need a target to belong to;
// this file is that target's only source.
