#include "gl/resource/query.h"

#include "gl/debug.h"
#include "gl/gl.h"

namespace bounce::gl {

void QueryDeleter::operator()(unsigned id) const
{
    glDeleteQueries(1, &id);
}

namespace {

// GL_ARB_pipeline_statistics_query's targets: Mesa's glCreateQueries refuses them (GL_INVALID_ENUM), so
// their names come from glGenQueries and exist as objects from their first glBeginQuery.
bool isPipelineStatistic(unsigned target)
{
    return (target >= 0x82EE && target <= 0x82F7) || target == 0x82F9 || target == 0x8F9B || target == 0x82F2;
}

} // namespace

Query::Query(unsigned target, const std::string& label) : target_(target)
{
    unsigned id = 0;
    if (isPipelineStatistic(target)) {
        glGenQueries(1, &id);
        label_ = label; // labelled at the first begin(), when the object exists
    } else {
        glCreateQueries(target, 1, &id);
        labelObject(GL_QUERY, id, label);
    }
    handle_ = Handle<QueryDeleter>(id);
}

void Query::begin()
{
    if (!handle_) throw QueryError("begin on an empty query");
    if (active_) throw QueryError("begin on a query that is already active");
    glBeginQuery(target_, handle_.id());
    if (!label_.empty()) {
        labelObject(GL_QUERY, handle_.id(), label_);
        label_.clear();
    }
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
