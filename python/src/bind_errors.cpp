// tandem.Error: what the library's Status and Result errors become in Python; tandem.IdError:
// the same for an id the world does not hold.
#include "bindings.h"

namespace tandem::python {

void bindErrors(py::module_& module) {
  static py::exception<LibraryError> error(module, "Error", PyExc_RuntimeError);
  error.doc() =
      "An error the Tandem library reported (bad input refused, a step that diverged, a scene "
      "file that does not load). str(e) is the library's message, e.g. "
      "'rope: node count must be >= 2, got 1'.";
  // Both a tandem.Error and an IndexError: `except tandem.Error` and `except IndexError` both catch it.
  static py::exception<IdError> idError(module, "IdError", py::make_tuple(error, py::handle(PyExc_IndexError)));
  idError.doc() =
      "An id the world does not hold: never made, or stale (what it named was removed; its slot may "
      "hold something newer). A tandem.Error and an IndexError; str(e) names the call and the id, e.g. "
      "'rigid_position: rigid body 2 (generation 0) was removed'.";
  py::register_exception_translator([](std::exception_ptr pending) {
    try {
      if (pending) std::rethrow_exception(pending);
    } catch (const IdError& e) {
      idError(e.what());
    } catch (const LibraryError& e) {
      error(e.what());
    }
  });
}

}  // namespace tandem::python
