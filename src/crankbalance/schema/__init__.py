"""The descriptions of crankbalance's inputs: the engine file (:mod:`.engine`) and the
settings of every study (:mod:`.settings`), both declared with the machinery of
:mod:`.core`, from which validation, the documentation's tables and a JSON Schema are
derived."""
