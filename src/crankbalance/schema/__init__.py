"""The descriptions of crankbalance's inputs: the engine file (:mod:`.engine`) and the
settings of every study (:mod:`.settings`)."""
