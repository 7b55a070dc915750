"""The study layer: every derivation from an engine (file, preset, spec or model) to the
input of a physics study, and the orchestration of a whole study.

The command line, the web application and the report call this layer and nothing below
it for engine-derived quantities, so that one question has one answer everywhere:

* :mod:`.build`: engine spec -> :class:`~crankbalance.physics.model.EngineModel` (SI arrays).
* :mod:`.engine`: free forces and moments (:func:`.engine.analyze`) and the
  counterweights and balance shafts (:func:`.engine.balance_engine`).
* :mod:`.cylinder`: one cylinder of an engine (the shared-crankpin rule), its
  balance-factor study, the ISO 21940-11 check and its rebalancing.
* :mod:`.requirements`: the first moment a crank counterweight and the unbalance a
  balance shaft must carry, from the balancing solver.
* :mod:`.performance`: one cylinder as the engine-cycle model sees it.
"""
