// ref/ placeholder translation unit (replaced by the path tracer)
