"""The contact law in scaled units: internal scales, the MDR law, its branches and cascades,
spring arrays, the Maugis–Dugdale law."""
