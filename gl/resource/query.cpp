#include "gl/resource/query.h"

#include "gl/debug.h"
#include "gl/gl.h"

namespace bounce::gl {

void QueryDeleter::operator()(unsigned id) const
{
    glDeleteQueries(1, &id);
}

Query::Query(unsigned target, const std::string& label) : target_(target)
{
    unsigned id = 0;
    glCreateQueries(target, 1, &id);
    handle_ = Handle<QueryDeleter>(id);
    labelObject(GL_QUERY, id, label);
}

void Query::begin()
{
    if (!handle_) throw QueryError("begin on an empty query");
    if (active_) throw QueryError("begin on a query that is already active");
    glBeginQuery(target_, handle_.id());
    active_ = true;
}

void Query::end()
{
    if (!active_) throw QueryError("end on a query that is not active");
    glEndQuery(target_);
    active_ = false;
    ended_ = true;
}

Query::Scope Query::scope()
{
    begin();
    return Scope(this);
}

bool Query::resultAvailable() const
{
    if (!ended_ || active_) return false;
    GLuint available = GL_FALSE;
    glGetQueryObjectuiv(handle_.id(), GL_QUERY_RESULT_AVAILABLE, &available);
    return available == GL_TRUE;
}

std::uint64_t Query::result() const
{
    if (!ended_ || active_) throw QueryError("result of a query that has not ended");
    GLuint64 value = 0;
    glGetQueryObjectui64v(handle_.id(), GL_QUERY_RESULT, &value);
    return value;
}

} // namespace bounce::gl
