"""The validation and robustness suites (docs/validation.md, docs/stability.md) and the thesis's
chapter 5 (docs/thesis-figures.md), each a command of the package."""
