"""The descriptions of every input of crankbalance: the engine file, the settings of every
study, and the machinery (:mod:`.core`) from which validation, command-line options, the web
form, the documentation's tables and a JSON Schema are derived."""
