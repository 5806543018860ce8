#pragma once
// A reference to something callable with its type left out, like C++26's std::function_ref: it
// owns nothing, so the callable must outlive it. It lets a loop that is compiled once, in
// zraka::compiled (compiled.hpp), call a program's own lambda: one call through a pointer each
// time, instead of compiling the loop again for every lambda of every program. It refers to an
// object (a lambda, a functor); wrap a plain function in a lambda.
#include <memory>
#include <type_traits>
#include <utility>

namespace zraka {

template <class Signature> class function_ref;

template <class R, class... Args> class function_ref<R(Args...)> {
 public:
  template <class F>
    requires(!std::is_same_v<std::remove_cvref_t<F>, function_ref> && !std::is_function_v<std::remove_reference_t<F>> &&
             std::is_invocable_v<F&, Args...>)
  function_ref(F&& f)  // implicit, so that a lambda is passed as it is
      : obj_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
        call_([](void* o, Args... a) -> R {
          return R((*static_cast<std::remove_reference_t<F>*>(o))(std::forward<Args>(a)...));
        }) {}

  R operator()(Args... a) const { return call_(obj_, std::forward<Args>(a)...); }

 private:
  void* obj_;
  R (*call_)(void*, Args...);
};

}  // namespace zraka
