"""Output edges: formatting of numbers and units for people (:mod:`.format`), figures
(:mod:`.figures`), rendering to PNG, SVG, HTML and PDF (:mod:`.render`), reports
(:mod:`.report`) and the balance shop sheet (:mod:`.shop_sheet`)."""
