"""The post-processor example of python/README.md, run as written: its
```python blocks are executed and every `test_` function they define is
called."""

import pathlib
import re

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def blocks():
    return re.findall(r"```python\n(.*?)```", README.read_text(), re.S)


def test_the_readme_example_runs_and_passes():
    example = [b for b in blocks() if "def test_" in b]
    assert example, "the README lost its post-processor example"
    namespace = {}
    exec(compile("\n".join(example), str(README), "exec"), namespace)
    tests = [f for name, f in namespace.items() if name.startswith("test_")]
    assert len(tests) == 2
    for t in tests:
        t()
