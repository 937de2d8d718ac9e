// SPDX-License-Identifier: LGPL-3.0-or-later
// Empty: the target that compiles the precompiled headers (see CMakeLists.txt).
