# The extension module (python/bindings/): an internal interface, typed through the package's modules.
from typing import Any

def __getattr__(name: str) -> Any: ...
