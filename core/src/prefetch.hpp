// Asking memory for data ahead of its use, in a form the optimiser cannot drop.
#pragma once

#include <cstdint>

namespace softstep {

// Starts loading the cache line that holds `address` into every cache level (prefetcht0 on
// x86). Not __builtin_prefetch: gcc 12 deletes it where it judges it to have no effect. Its
// pure-const pass finds a function made only of prefetches `const`, and a call to a const
// function that returns nothing is dropped; a loop made only of prefetches is deleted as a
// finite loop without side effects (-ffinite-loops, on from -O2 in C++11 and later). The
// contacts' packing pass lost every prefetch that way without a word (`objdump -d`: none).
// A volatile asm is never removed. Both kinds of access use the read hint: prefetchw is not
// part of the portable build's instruction set.
inline void prefetch_line(const void* address) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(address)));
#else
  __builtin_prefetch(address);
#endif
}

// Every cache line the object touches (an object that does not start on a line's start
// reaches into one more line than sizeof / 64).
template <class T>
void prefetch_object(const T& object) {
  const auto begin = reinterpret_cast<std::uintptr_t>(&object) & ~std::uintptr_t{63};
  const auto end = reinterpret_cast<std::uintptr_t>(&object) + sizeof(T);
  for (std::uintptr_t at = begin; at < end; at += 64)
    prefetch_line(reinterpret_cast<const void*>(at));
}

}  // namespace softstep
