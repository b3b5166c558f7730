// gl/ placeholder translation unit
