// Reading a glTF file's data back in tests: an accessor's values as a flat array.
#pragma once
#include <cstring>
#include <vector>

#include <tiny_gltf.h>

namespace lrigid::test {

// accessor `index` of `m` as count x comps values of T (tightly packed, as the writers lay them)
template <typename T>
std::vector<T> accessor_data(const tinygltf::Model& m, int index, int comps) {
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
  const unsigned char* p = m.buffers[size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  std::vector<T> out(a.count * size_t(comps));
  std::memcpy(out.data(), p, out.size() * sizeof(T));
  return out;
}

}  // namespace lrigid::test
