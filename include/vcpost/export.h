// What the shared library libvcpost exports: the classes and functions of
// <vcpost/...> only. Everything else in it is internal and hidden, so the
// internals can change without breaking a program linked against it.
#pragma once

#define VCPOST_API __attribute__((visibility("default")))
